// gazebo_plugins' publishing queues (car's drop-in; behaviour of gazebo_ros_pkgs noetic-devel
// gazebo_plugins/include/gazebo_plugins/PubQueue.h, written for car): a plug-in pushes (message, publisher) pairs
// from the physics thread onto a PubQueue<T>; a PubMultiQueue's service thread publishes every pair pushed, in the
// order pushed, so the physics thread does not wait on ROS. Unlike upstream's, a push made while the thread is busy
// is never left waiting for the next push.
#pragma once

#include <boost/bind.hpp>
#include <boost/function.hpp>
#include <boost/shared_ptr.hpp>
#include <boost/thread.hpp>
#include <deque>
#include <list>
#include <ros/ros.h>
#include <vector>

// One message and the publisher it goes out on.
template <class T>
class PubMessagePair {
 public:
  T msg_;
  ros::Publisher pub_;
  PubMessagePair(T& msg, ros::Publisher& pub) : msg_(msg), pub_(pub) {}
};

// The pairs of one message type waiting for the service thread.
template <class T>
class PubQueue {
 public:
  typedef boost::shared_ptr<std::deque<boost::shared_ptr<PubMessagePair<T> > > > QueuePtr;
  typedef boost::shared_ptr<PubQueue<T> > Ptr;

  PubQueue(QueuePtr queue, boost::shared_ptr<boost::mutex> queue_lock, boost::function<void()> notify_func)
      : queue_(queue), queue_lock_(queue_lock), notify_func_(notify_func) {}

  // Copies the message and wakes the service thread.
  void push(T& msg, ros::Publisher& pub) {
    boost::shared_ptr<PubMessagePair<T> > pair(new PubMessagePair<T>(msg, pub));
    {
      boost::mutex::scoped_lock lock(*queue_lock_);
      queue_->push_back(pair);
    }
    notify_func_();
  }

  // Moves every waiting pair to the end of els, oldest first.
  void pop(std::vector<boost::shared_ptr<PubMessagePair<T> > >& els) {
    boost::mutex::scoped_lock lock(*queue_lock_);
    els.insert(els.end(), queue_->begin(), queue_->end());
    queue_->clear();
  }

 private:
  QueuePtr queue_;
  boost::shared_ptr<boost::mutex> queue_lock_;
  boost::function<void()> notify_func_;
};

// The queues of a plug-in and the thread that publishes what they hold.
class PubMultiQueue {
 public:
  PubMultiQueue() {}
  ~PubMultiQueue() {
    {
      boost::mutex::scoped_lock lock(wake_lock_);
      running_ = false;
      ++pending_;
    }
    wake_.notify_one();
    if (thread_.joinable()) thread_.join();
  }

  // A new queue for messages of type T, served by this object.
  template <class T>
  boost::shared_ptr<PubQueue<T> > addPub() {
    typename PubQueue<T>::QueuePtr queue(new std::deque<boost::shared_ptr<PubMessagePair<T> > >);
    boost::shared_ptr<boost::mutex> lock(new boost::mutex);
    boost::shared_ptr<PubQueue<T> > pq(new PubQueue<T>(queue, lock, boost::bind(&PubMultiQueue::notifyServiceThread, this)));
    boost::mutex::scoped_lock funcs(funcs_lock_);
    funcs_.push_back(boost::bind(&PubMultiQueue::publishAll<T>, this, pq));
    return pq;
  }

  // Publishes what every queue holds now, on the calling thread.
  void spinOnce() {
    boost::mutex::scoped_lock lock(funcs_lock_);
    for (auto& f : funcs_) f();
  }

  // Publishes as pushes come, until ROS shuts down or this object goes.
  void spin() {
    while (ros::ok()) {
      {
        boost::unique_lock<boost::mutex> lock(wake_lock_);
        while (pending_ == 0) wake_.wait(lock);
        pending_ = 0;
        if (!running_) return;
      }
      spinOnce();
    }
  }

  void startServiceThread() {
    {
      boost::mutex::scoped_lock lock(wake_lock_);
      running_ = true;
    }
    thread_ = boost::thread(boost::bind(&PubMultiQueue::spin, this));
  }

  void notifyServiceThread() {
    {
      boost::mutex::scoped_lock lock(wake_lock_);
      ++pending_;
    }
    wake_.notify_one();
  }

 private:
  template <class T>
  void publishAll(boost::shared_ptr<PubQueue<T> > pq) {
    std::vector<boost::shared_ptr<PubMessagePair<T> > > els;
    pq->pop(els);
    for (auto& el : els) el->pub_.publish(el->msg_);
  }

  std::list<boost::function<void()> > funcs_;
  boost::mutex funcs_lock_;
  boost::thread thread_;
  boost::mutex wake_lock_;
  boost::condition_variable wake_;
  unsigned pending_ = 0;
  bool running_ = false;
};
